"""The examples that ship with the package, so that every snippet of the site runs from any folder
after ``pip install uwml``: robot descriptions with their hydro files, logs and study files
(:func:`path`, :func:`bluerov2`, :func:`my_arm`), and a robot made in code (:func:`arm_on_rov`).
Their numbers are illustrative where they are not a vehicle's published ones (each file says).

======================  =====================================================================
``path(...)``           what
======================  =====================================================================
``"bluerov2"``          a BlueROV2 Heavy with a 2-joint arm: ``bluerov2_arm.urdf``, its hydro
                        file ``bluerov2_arm.hydro.toml`` (Fossen's lumped hull with published
                        parameters, eight thrusters), a free-running log ``dive.csv`` and the
                        script that made it, a README
``"my_arm"``            a 2-joint arm: ``my_arm.urdf``, ``my_arm.hydro.toml``, a land/water
                        log ``land_water.csv``, a water-only log ``water.csv``, and the
                        scripts that made them
``"mjx_rollout.py"``    a batched rollout of the BlueROV2 in MJX with a reward (``uwml[jax]``)
``"hydro.toml"``        a hydro file showing every key
``"study.toml"``        a study of the paper's leg; ``"vehicle_study.toml"`` one of the
                        BlueROV2 keeping station
======================  =====================================================================
"""

from .code_robots import arm_on_rov
from .shipped import bluerov2, my_arm, names, path

__all__ = ["arm_on_rov", "bluerov2", "my_arm", "names", "path"]
