"""The command line the A/B benches share: ``--base`` (a folder holding the
other build, importable as ``splinelab_base``), ``--rounds`` and the case
names; returns the arguments and the two builds, ours and the base."""

import argparse
import sys


def parse_ab(rounds=7):
    """``(args, splinelab, splinelab_base)`` from ``sys.argv``."""
    p = argparse.ArgumentParser()
    p.add_argument("--base", required=True, help="folder holding the other build as splinelab_base")
    p.add_argument("--rounds", type=int, default=rounds)
    p.add_argument("cases", nargs="*")
    args = p.parse_args()
    sys.path.insert(0, args.base)
    import splinelab
    import splinelab_base

    return args, splinelab, splinelab_base
