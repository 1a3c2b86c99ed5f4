"""The engine of the GLD fits: compiled shape equations and objectives, their solvers, the
candidate solutions and the sample statistics they match (no public names; the public fits are
in :mod:`glstat.fitting`)."""
