"""bearing_core: angular-contact ball bearing models (Hertz contact, Jones-Harris quasi-statics, pure
rolling lines, Gupta-style tribo-dynamics in numba). SI units inside; see README.md."""
