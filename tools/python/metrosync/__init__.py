"""metrosync from Python: coupled metronomes on a platform with dry friction.

    import metrosync
    res = metrosync.run("yaml/rigs/experiment.yaml", duration=60)    # a path, a dict or a Rig
    res.regime, res.envelope["A_1"], res.to_pandas()                 # numpy arrays, a DataFrame
    rig = metrosync.load_rig("yaml/rigs/experiment.yaml", {"platform.friction.mu": 0.3})
    grid = metrosync.sweep(rig, vary={"platform.friction.mu": (0, 1, 21)})
    grid.regime, grid["A_1"]                                         # arrays shaped by the grid

Every call runs the command-line program's own code in-process (the same C++ functions), its
rows kept in memory: the arrays hold the numbers the CLI's files print (to 12 digits). Files are
written only into ``out=DIR``. docs/python.md is the reference.
"""

from . import _metrosync as _core
from ._calls import basin, compare, continue_, fit, run, sweep
from ._results import (BasinResult, CompareResult, ContinuationResult, FitResult, Result,
                       SimulationError, SweepResult)
from ._rig import Rig, RigError, load_rig

__all__ = ["Rig", "Result", "CompareResult", "SweepResult", "BasinResult", "ContinuationResult",
           "FitResult", "RigError", "SimulationError", "load_rig", "run", "compare", "sweep",
           "basin", "continue_", "fit", "version"]


def version():
    """metrosync's version (as ``metrosync --version`` prints it first).

    >>> metrosync.version()
    '0.1.0'
    """
    return _core.version()
