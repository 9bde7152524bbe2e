"""Bearing models: Jones-Harris quasi-statics (two- and four-point contact), the tribological quasi-static
model, the Gupta-style dynamics (kernels, integrators, Python API), skid classification and wear."""
