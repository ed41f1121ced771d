"""What a robot is made of, as plain checked numbers: its parts (:mod:`uwml.model.parts`: joints,
links, segments, the water), its joints' losses (:mod:`uwml.model.losses`: drive, oil drag,
seal; :mod:`uwml.model.joint_losses`: a joint's losses together, evaluated by the Rust core) and
lumped hydrodynamic models (:mod:`uwml.model.lumped`).

The package imports only the pure-Python :mod:`~uwml.model.parts` and :mod:`~uwml.model.losses`;
:mod:`uwml.model.joint_losses` (which needs the compiled core) and :mod:`uwml.model.lumped` are
imported when named.
"""

from .losses import Drive, OilDrag, Seal
from .parts import (
    CIRCULAR_DEFAULTS,
    FRESH_WATER,
    RECTANGULAR_DEFAULTS,
    SEA_WATER,
    SECTIONS,
    Joint,
    Link,
    Segment,
    Vec3,
    Water,
)

__all__ = [
    "CIRCULAR_DEFAULTS",
    "FRESH_WATER",
    "RECTANGULAR_DEFAULTS",
    "SEA_WATER",
    "SECTIONS",
    "Drive",
    "Joint",
    "Link",
    "OilDrag",
    "Seal",
    "Segment",
    "Vec3",
    "Water",
]
