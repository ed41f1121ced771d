"""The sea around a joint: depth, pressure and temperature (:mod:`uwml.sea.conditions`), sea water
by TEOS-10 (:mod:`uwml.sea.seawater`) and the compensation oil's viscosity (:mod:`uwml.sea.oil`).

Pure Python and numpy (``gsw`` for TEOS-10): no compiled code. The package imports only
:mod:`~uwml.sea.conditions`; the other two are imported when named.
"""

from .conditions import (
    ExtrapolationWarning,
    check_depths,
    check_temperatures,
    hydrostatic_pressure,
    hydrostatic_pressure_mpa,
    positive_number,
)

__all__ = [
    "ExtrapolationWarning",
    "check_depths",
    "check_temperatures",
    "hydrostatic_pressure",
    "hydrostatic_pressure_mpa",
    "positive_number",
]
