"""whirl: the physics of a chain spun about the vertical axis, from Python (numpy arrays over the
C library libwhirl, through cffi).

Steady shapes: critical, shape, sweep, equilibria. Dynamics: Chain, Simulation. Stability:
stability, stability_map, stability_windows, dissipative_windows, atlas. The hand-swung chain:
driven, driven_branch, spin_up. Measured shapes: fit. Scene files: run_scene. whirl's CSV
files: read_csv.
A pivot on a periodic path: periodic (a periodic motion and its Floquet multipliers),
periodic_path (a branch of them), chart_vertical (the shaken chain's stability chart),
chart_ellipse (the hand-swung chain's ellipticity chart).
Units follow the command line's rule (whirl.Units): dimensionless (chain length, mass and
gravity = 1) unless length [m], mass [kg] or gravity [m/s^2] is given, or a Units object; then
SI, gravity defaulting to 9.80665 m/s^2. Library failures raise whirl.Error with the library's
message (bad values: whirl.InvalidInput, also a ValueError); Ctrl-C during a long call raises
KeyboardInterrupt naming the call; the calls that can take seconds take progress= (None; True:
a tqdm bar, or a line on standard error; or a callable (done, total)). Results are dataclasses
that pickle and copy; as_dict() and to_pandas() give their tables in the command line's column
names with units (whirl.columns). Numbers with a unit may be texts ("4Hz") or pint quantities;
shape() over an array of rates returns Shapes. A run whose fixed step damping or drag makes stiff
takes gsl-msbdf with a StiffWarning unless its method was named.
Threads: a Simulation serves one thread at a time (a second thread gets whirl.InUse); the
library's own parallel loops take whirl.max_threads() OpenMP threads (whirl.set_max_threads),
one in a child of fork().
``whirl.__version__`` is the library's version; ``whirl.LIBRARY_PATH`` the library in use."""
from ._lib import (Error, InUse, InvalidInput, LIBRARY_PATH, LIBRARY_VERSION, max_threads,
                   methods, set_max_threads, stop_requested)
from .steady import (STANDARD_GRAVITY, EmptyBranchWarning, Units, Chain, Shape, Shapes, critical,
                     equilibria, shape, sweep)
from .dynamics import Simulation, StiffWarning, Trajectory
from .stability import (StabilityResult, dissipative_windows, stability, stability_map,
                        stability_windows)
from .driven import DrivenShape, SpinUp, driven, spin_up
from .driven import DrivenBranch, driven_branch
from .atlas import atlas
from .fit import FitResult, fit
from .scene import SceneRun, run_scene
from .csv import Table, read_csv
from .periodic import (Chart, EllipseChart, PeriodicBranch, PeriodicResult, chart_ellipse,
                       chart_vertical, periodic, periodic_path)

__version__ = LIBRARY_VERSION

__all__ = ["Error", "InUse", "InvalidInput", "LIBRARY_PATH", "methods", "stop_requested",
           "max_threads", "set_max_threads",
           "STANDARD_GRAVITY", "EmptyBranchWarning", "Units", "Chain", "Shape", "Shapes", "critical",
           "equilibria", "shape",
           "sweep", "Simulation", "StiffWarning", "Trajectory", "StabilityResult", "stability",
           "stability_map", "stability_windows", "dissipative_windows", "DrivenShape", "SpinUp",
           "driven", "spin_up",
           "DrivenBranch", "driven_branch", "atlas",
           "FitResult", "fit", "SceneRun", "run_scene", "Table", "read_csv",
           "PeriodicResult", "PeriodicBranch", "Chart", "periodic", "periodic_path",
           "chart_vertical", "EllipseChart", "chart_ellipse", "__version__"]
