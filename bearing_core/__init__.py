"""bearing_core: angular-contact ball bearing models (Hertz contact, Jones-Harris quasi-statics, pure
rolling lines, Gupta-style tribo-dynamics in numba). SI units inside; see README.md."""
# scipy's Fortran runtime is loaded before numba/llvmlite on purpose: the reverse order made processes that
# host the bearing FMU abort at exit with heap corruption (docs/fmu.md).
import scipy.linalg  # noqa: F401
