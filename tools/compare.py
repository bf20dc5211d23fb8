#!/usr/bin/python3
"""Compare an impact3d dump with the exact solution of a verification problem:
the command line of impact3d_tools.compare (its docstring defines the
problems, norms and shock measures; --help lists the options).

Usage: tools/compare.py --problem {sod,riemann2,sedov,noh} dump.h5 [--out summary.txt] ...
"""
import sys

from impact3d_tools import compare

if __name__ == "__main__":
    sys.exit(compare.main())
