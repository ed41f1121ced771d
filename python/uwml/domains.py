"""The domains of the physics' inputs (docs/domains.md), in pure Python so that the modules that
need no compiled core (``seawater``, ``oil``, ...) can check them too. The Rust core holds the
same numbers (``uwml_core::MAX_DEPTH`` and the others); a test holds the two equal."""

#: The deepest ocean [m]: depths are taken from 0 to this (the Challenger Deep is about 10,935 m).
MAX_DEPTH = 11_000.0
#: The largest ambient (gauge) pressure taken [Pa]: the deepest ocean's 110 MPa, with margin.
MAX_PRESSURE = 1.2e8
#: The most joints of a robot built from Python (``uwml.MAX_ROBOT_JOINTS``), and so of a log.
MAX_ROBOT_JOINTS = 64
#: Absolute zero [°C]: temperatures must be above it.
ABSOLUTE_ZERO_C = -273.15
#: The oil temperatures [°C] the oil model is meant for: the sea's, from where sea water freezes
#: (about −2 °C) to the 40 °C of the oil's viscosity grade.
OIL_TEMPERATURE_RANGE_C = (-2.0, 40.0)

# A model's values (docs/domains.md, "Model values"): larger is a unit mistake, or a value whose
# forces would overflow. Every coordinate of a point and every length, width and diameter [m]:
MAX_LENGTH = 1e4
#: A body's mass [kg] (the largest ships displace under 1e9 kg).
MAX_MASS = 1e9
#: A body's volume [m³].
MAX_VOLUME = 1e6
#: A segment's cross-section area [m²].
MAX_AREA = 1e8
#: A drag or added-mass coefficient (measured ones are of order 1).
MAX_COEFFICIENT = 1e3
#: A water's density [kg/m³] (more than any liquid's).
MAX_DENSITY = 1e5
#: Gravity [m/s²].
MAX_GRAVITY = 1e3
