"""Contact mechanics: Hertz point contact and its tables, Jones-Harris ball kinematics, pure-rolling lines and
spin friction, Kalker's FASTSIM, the traction-parameter layout and per-contact numba kernels."""
