"""The `trnkit` command of a pip install (pyproject.toml's console script): runs the CLI that the
wheel carries as trnkit/bin/trnkit (built from apps/trnkit with the package's own libraries), with
the same arguments, exit status and output as `trnkit` from a CMake build."""
import os
import sys


def executable():
    """The CLI beside this package, or None (a package assembled by the CMake build, not by pip: there
    the CLI is build/apps/trnkit/trnkit, and `cmake --install` puts it in bin/)."""
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bin", "trnkit")
    return path if os.access(path, os.X_OK) else None


def main():
    path = executable()
    if path is None:
        sys.stderr.write("trnkit: this trnkit package has no CLI (trnkit/bin/trnkit): it comes with `pip install`; a CMake "
                         "build has it as build/apps/trnkit/trnkit\n")
        return 2
    os.execv(path, ["trnkit", *sys.argv[1:]])
    return 0  # not reached


if __name__ == "__main__":
    sys.exit(main())
