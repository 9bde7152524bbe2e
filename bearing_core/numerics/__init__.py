"""Numerics shared by every layer: compile flags of the hot kernels (jit) and error-bounded polynomial
elementary functions (mathx)."""
