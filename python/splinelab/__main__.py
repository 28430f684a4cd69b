"""``python -m splinelab`` and the wheel's ``splinelab`` console script.

The same command line as the Rust binary (``splinelab check``, ``compare``,
``report``, ...), run by the extension, so ``pip install splinelab`` gives
it without a Rust toolchain. Exit statuses as the binary's (``--help``).
"""

from __future__ import annotations

import sys


def main(argv: list[str] | None = None) -> int:
    """Run ``splinelab ARGS`` and return its exit status.

    Parameters
    ----------
    argv : list of str, optional
        The arguments after ``splinelab`` (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        The exit status, as the Rust binary's (``splinelab --help``).

    Examples
    --------
    >>> from splinelab.__main__ import main
    >>> main(["--version"])  # doctest: +ELLIPSIS
    splinelab ...
    0
    """
    from . import _splinelab as _ext

    args = sys.argv[1:] if argv is None else list(argv)
    # The command prints through the process's own stdout: what Python
    # buffered so far goes first.
    sys.stdout.flush()
    sys.stderr.flush()
    return _ext.cli_main(["splinelab", *args])


if __name__ == "__main__":
    sys.exit(main())
