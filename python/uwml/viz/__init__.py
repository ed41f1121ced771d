"""What a person looks at: figures of the joint losses and of the fits (:mod:`uwml.viz.plot`,
matplotlib) and a robot described in words and drawn (:mod:`uwml.viz.describe`).

The package imports none of its modules (matplotlib is imported with :mod:`uwml.viz.plot`).
"""
