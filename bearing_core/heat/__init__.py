"""Heat: the bearing's thermal network (nodes, conductances, steady and transient solves, runaway)."""
