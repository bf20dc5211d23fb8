#!/usr/bin/python3
"""Plot zone profiles of an impact3d dump against the exact solution: the
command line of impact3d_tools.profiles (--help lists the options).

Usage: tools/plot_profiles.py --problem {sod,riemann2,sedov,noh} dump.h5 [-o out.png] ...
"""
import sys

from impact3d_tools import profiles

if __name__ == "__main__":
    sys.exit(profiles.main())
