"""Run by capi.installed_consumers with PYTHONPATH at an installed prefix (argv[1]): the module
found is the installed one, and it loads libtrnkit through its RUNPATH (gx of a ramp rising 10 per
column: 4 x 20 = 80)."""
import sys

import numpy as np

import trnkit

assert trnkit.__file__.startswith(sys.argv[1]), trnkit.__file__
gx, gy = trnkit.Backend("cpu").sobel(np.tile(np.arange(0, 80, 10, dtype=np.uint8), (8, 1)))
print("python: installed trnkit", trnkit.__version__, "gx", int(gx[3, 3]))
