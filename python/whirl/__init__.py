"""whirl: the physics of a chain spun about the vertical axis, from Python (numpy arrays over the
C library libwhirl, through cffi).

Steady shapes: critical, shape, sweep, equilibria. Dynamics: Chain, Simulation. Stability:
stability, stability_map, stability_windows. The hand-swung chain: driven, spin_up. Measured
shapes: fit. Scene files: run_scene.
Units are dimensionless (chain length, mass and gravity = 1) unless length [m], mass [kg] and
gravity [m/s^2] are given. Library failures raise whirl.Error with the library's message;
Ctrl-C during a long call raises KeyboardInterrupt."""
from ._lib import Error, LIBRARY_PATH, methods, stop_requested
from .steady import Units, Chain, Shape, critical, equilibria, shape, sweep
from .dynamics import Simulation, Trajectory
from .stability import StabilityResult, stability, stability_map, stability_windows
from .driven import DrivenShape, SpinUp, driven, spin_up
from .fit import FitResult, fit
from .scene import SceneRun, run_scene

__all__ = ["Error", "LIBRARY_PATH", "methods", "stop_requested", "Units", "Chain", "Shape",
           "critical", "equilibria", "shape", "sweep", "Simulation", "Trajectory",
           "StabilityResult",
           "stability", "stability_map", "stability_windows", "DrivenShape", "SpinUp", "driven", "spin_up",
           "FitResult", "fit", "SceneRun", "run_scene"]
