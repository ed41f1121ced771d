"""What a robot is made of, as plain checked numbers: its parts (:mod:`uwml.model.parts`: joints,
links, segments, the water) and its joints' losses (:mod:`uwml.model.losses`: drive, oil drag,
seal; :mod:`uwml.model.joint_losses`: a joint's losses together, evaluated by the Rust core).

The package imports only the pure-Python :mod:`~uwml.model.parts` and :mod:`~uwml.model.losses`
(it keeps the names of the former module ``uwml.model``); :mod:`uwml.model.joint_losses`, which
needs the compiled core, is imported when named.
"""

from .._checks import to_float as to_float
from ..domains import MAX_DENSITY as MAX_DENSITY
from ..domains import MAX_GRAVITY as MAX_GRAVITY
from .losses import RPM as RPM
from .losses import Drive as Drive
from .losses import OilDrag as OilDrag
from .losses import Seal as Seal
from .parts import AXIS_TOLERANCE as AXIS_TOLERANCE
from .parts import CIRCULAR_DEFAULTS, RECTANGULAR_DEFAULTS, SECTIONS, Joint, Link, Segment, Vec3, Water
from .parts import FRESH_WATER as FRESH_WATER
from .parts import JOINT_KINDS as JOINT_KINDS
from .parts import SEA_WATER as SEA_WATER

__all__ = ["CIRCULAR_DEFAULTS", "RECTANGULAR_DEFAULTS", "SECTIONS", "Joint", "Link", "Segment", "Vec3", "Water"]
