"""A stand-in for sewar (https://github.com/andrewekhalel/sewar), which Debian does not package.

The 3D Commerce suite's evaluation.py imports vifp and uqi from it but never calls them (their
lines in evaluate_metrics are commented out), so these are never reached; they fail loudly if a
later evaluation.py starts to use them.
"""


def vifp(*_args, **_kwargs):
    raise NotImplementedError("sewar is not installed: scripts/certify/sewar stands in for its import only")


def uqi(*_args, **_kwargs):
    raise NotImplementedError("sewar is not installed: scripts/certify/sewar stands in for its import only")
