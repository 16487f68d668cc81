"""The argparse parser of every command: usage errors printed escaped (text.shown)."""
from __future__ import annotations

import argparse
import sys

from ..io import InputError
from ..text import shown


class Parser(argparse.ArgumentParser):
    """argparse's parser whose usage errors (which quote the offending argument) are
    printed escaped; subparsers inherit it."""

    def error(self, message: str):
        super().error(shown(message))


def fail(path: str, err: InputError) -> int:
    where = f"{path}:{err.where}" if err.where else path
    print(f"sva-tools: error: {shown(where)}: {shown(err)}", file=sys.stderr)
    return 2
