#!/usr/bin/python3
"""Entry point of the regression checks (package checks/, one module per kind
of check): check.py SUBCOMMAND --exe EXE --workdir DIR --deck DECK ...;
check.py --help lists the subcommands. Needs tools/ on PYTHONPATH."""
import sys

from checks import main

sys.exit(main())
