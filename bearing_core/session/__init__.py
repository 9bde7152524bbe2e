"""The FMI-free co-simulation session: inputs held over a step, rollback state, outputs as one array."""
