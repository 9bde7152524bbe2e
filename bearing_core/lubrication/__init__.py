"""Lubrication: oils and their rheology, Hamrock-Dowson film thickness, EHL traction over the Hertz ellipse,
the lubricated ball-pocket contact, churning, and the SKF 2004 / Palmgren friction estimates."""
