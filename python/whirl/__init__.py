"""whirl: the physics of a chain spun about the vertical axis, from Python (numpy arrays over the
C library libwhirl, through cffi).

Steady shapes: critical, shape, sweep, equilibria. Dynamics: Chain, Simulation. Stability:
stability, stability_map, stability_windows, dissipative_windows. The hand-swung chain: driven, spin_up. Measured
shapes: fit. Scene files: run_scene. whirl's CSV files: read_csv.
A pivot on a periodic path: periodic (a periodic motion and its Floquet multipliers),
periodic_path (a branch of them), chart_vertical (the shaken chain's stability chart).
Units follow the command line's rule (whirl.Units): dimensionless (chain length, mass and
gravity = 1) unless length [m], mass [kg] or gravity [m/s^2] is given, or a Units object; then
SI, gravity defaulting to 9.80665 m/s^2. Library failures raise whirl.Error with the library's
message (bad values: whirl.InvalidInput, also a ValueError); Ctrl-C during a long call raises
KeyboardInterrupt naming the call. Results are dataclasses that pickle and copy.
Threads: a Simulation serves one thread at a time (a second thread gets whirl.InUse); the
library's own parallel loops take whirl.max_threads() OpenMP threads (whirl.set_max_threads),
one in a child of fork().
``whirl.__version__`` is the library's version; ``whirl.LIBRARY_PATH`` the library in use."""
from ._lib import (Error, InUse, InvalidInput, LIBRARY_PATH, LIBRARY_VERSION, max_threads,
                   methods, set_max_threads, stop_requested)
from .steady import (STANDARD_GRAVITY, EmptyBranchWarning, Units, Chain, Shape, critical,
                     equilibria, shape, sweep)
from .dynamics import Simulation, Trajectory
from .stability import (StabilityResult, dissipative_windows, stability, stability_map,
                        stability_windows)
from .driven import DrivenShape, SpinUp, driven, spin_up
from .fit import FitResult, fit
from .scene import SceneRun, run_scene
from .csv import Table, read_csv
from .periodic import (Chart, PeriodicBranch, PeriodicResult, chart_vertical, periodic,
                       periodic_path)

__version__ = LIBRARY_VERSION

__all__ = ["Error", "InUse", "InvalidInput", "LIBRARY_PATH", "methods", "stop_requested",
           "max_threads", "set_max_threads",
           "STANDARD_GRAVITY", "EmptyBranchWarning", "Units", "Chain", "Shape", "critical",
           "equilibria", "shape",
           "sweep", "Simulation", "Trajectory", "StabilityResult", "stability",
           "stability_map", "stability_windows", "dissipative_windows", "DrivenShape", "SpinUp",
           "driven", "spin_up",
           "FitResult", "fit", "SceneRun", "run_scene", "Table", "read_csv",
           "PeriodicResult", "PeriodicBranch", "Chart", "periodic", "periodic_path",
           "chart_vertical", "__version__"]
