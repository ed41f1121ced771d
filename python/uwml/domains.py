"""The domains of the physics' inputs (docs/domains.md), in pure Python so that the modules that
need no compiled core (``seawater``, ``oil``, ...) can check them too. The Rust core holds the
same numbers (``uwml_core::MAX_DEPTH`` and the others); a test holds the two equal."""

#: The deepest ocean [m]: depths are taken from 0 to this (the Challenger Deep is about 10,935 m).
MAX_DEPTH = 11_000.0
#: The largest ambient (gauge) pressure taken [Pa]: the deepest ocean's 110 MPa, with margin.
MAX_PRESSURE = 1.2e8
#: Absolute zero [°C]: temperatures must be above it.
ABSOLUTE_ZERO_C = -273.15
#: The oil temperatures [°C] the oil model is meant for: the sea's, from where sea water freezes
#: (about −2 °C) to the 40 °C of the oil's viscosity grade.
OIL_TEMPERATURE_RANGE_C = (-2.0, 40.0)
