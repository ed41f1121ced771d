"""Files in and out: uwml model files (:mod:`uwml.io.modelfile`), robot descriptions URDF and
MJCF (:mod:`uwml.io.descriptions`) with their hydro files (:mod:`uwml.io.hydrofile`), C and Rust
source of a robot (:mod:`uwml.io.export`), and logs of joint states and torques
(:mod:`uwml.io.logs`, CSV and Parquet through pyarrow).

The readers give a robot's parts (joints, links, losses, water), which :mod:`uwml.robot`
assembles; the writers take any object with a robot's attributes. So io knows the model
(:mod:`uwml.model`), not the robots built on it. Every file is read only if it is a regular file
(a named pipe is refused, not waited on) and written whole or not at all.

The package imports none of its modules: name the one you need.
"""
