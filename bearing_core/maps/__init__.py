"""Operating maps: parameter sweeps of any model on Dask, with cache and resume."""
