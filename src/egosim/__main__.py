"""`python -m egosim` is the `egosim` command."""

from .cli import command

command()
