"""`python -I -S default_signals.py PROGRAM ARG...`: run PROGRAM with the signal handling a
program started from a shell has: no signal blocked, and SIGINT, SIGTERM, SIGPIPE and
SIGXFSZ at their default action.

A case's processes are started through it because a process inherits its parent's signal
mask and ignored signals across exec: Ray's workers block SIGINT, a shell's background job
ignores it, and Python ignores SIGPIPE and SIGXFSZ. Without it the SIGINT that stops a
case gracefully would never reach the case's simulator or stack on Ray. It imports only the
standard library (it runs without site-packages, in a few milliseconds).
"""

from __future__ import annotations

import os
import signal
import sys

RESET = (signal.SIGINT, signal.SIGTERM, signal.SIGPIPE, signal.SIGXFSZ)
EXIT_NOT_FOUND = 127
"""What a shell exits with for a command it cannot run."""


def main(argv: list[str]) -> int:
    if not argv:
        print("usage: default_signals.py PROGRAM [ARG...]", file=sys.stderr)
        return 2
    for number in RESET:
        signal.signal(number, signal.SIG_DFL)
    signal.pthread_sigmask(signal.SIG_SETMASK, ())
    try:
        os.execvp(argv[0], argv)
    except OSError as error:
        print(f"cannot run {argv[0]}: {error}", file=sys.stderr)
    return EXIT_NOT_FOUND


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
