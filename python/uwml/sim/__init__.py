"""Simulation of any robot: MuJoCo stepped with uwml's forces, the added mass in the mass matrix
(:mod:`uwml.sim.mujoco`, with the MJCF of a robot built in code, :mod:`uwml.sim.mjcf`), joint
motion prescribed or in closed form (:mod:`uwml.sim.prescribed`), a recorded arm motion replayed
on a floating vehicle (:mod:`uwml.sim.replay`, ``uwml replay``) and closed-loop control: tracking
and station keeping (:mod:`uwml.sim.control`; through a vehicle's thrusters, their curves
inverted: :mod:`uwml.sim.station_keeping`, :mod:`uwml.sim.thrust_inverse`). The paper's own
simulations are :mod:`uwml.paper`'s.

The package imports none of its modules: name the one you need (MuJoCo is imported when a
simulation is made).
"""
