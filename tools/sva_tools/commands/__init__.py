"""`sva-tools SUBCOMMAND ...`: one entry point for every host tool (docs/tools.md)."""
from __future__ import annotations

import importlib
import sys

from .. import __version__, io
from ..text import shown
from .common import Parser, fail

SUBCOMMANDS = ("gen", "check", "validate", "ref", "ih", "peer", "bench", "plot", "sim", "ground", "geo",
               "mavlink", "campaign", "sitl")


def _lcm(argv: list[str]) -> int:
    # `lcm` belongs to the LCM port's helper package sva_tools.lcm; it is
    # dispatched when present and reported clearly when not.
    try:
        mod = importlib.import_module("sva_tools.commands.lcm")
    except ImportError as e:
        print(f"sva-tools: error: the lcm subcommand is not available ({shown(e)}); it needs the "
              f"sva_tools.lcm package (LCM port) and the lcm Python module", file=sys.stderr)
        return 2
    return int(mod.main(argv))


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv and argv[0] == "lcm":
        return _lcm(argv[1:])
    ap = Parser(prog="sva-tools", description=__doc__)
    ap.add_argument("--version", action="version", version=f"sva-tools {__version__}",
                    help='print "sva-tools VERSION" (the sva library\'s) and exit')
    sub = ap.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    for name in SUBCOMMANDS:
        importlib.import_module(f"sva_tools.commands.{name}").add_parser(sub)
    sub.add_parser("lcm", help="LCM port tools (sva_tools.lcm, when installed)")
    args = ap.parse_args(argv)
    try:
        return int(args.func(args))
    except io.InputError as e:  # a bad mission or plan file (SPEC 4): one line, exit 2
        return fail(e.path or args.command, e)
    except KeyboardInterrupt:
        print(f"sva-tools: {args.command}: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        return 1

