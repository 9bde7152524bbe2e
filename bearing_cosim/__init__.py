"""Host-side tools for the bearing FMU: drive it with fmpy through speed/load profiles (the `bearing
simulate` command). Kept apart from bearing_core, which has no FMI knowledge."""
