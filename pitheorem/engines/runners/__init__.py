"""Runners: each compiles a format's document in its engine and runs it.

One module per engine, each with one line in
:data:`pitheorem.engines.registry.REGISTRY`: ``mujoco``, ``mjx`` (on
MuJoCo's compilation) and ``pybullet``.  A runner states its precision,
the numbers its engine stores, its options and remedies, and provides
what :mod:`pitheorem.engines.protocols` names; only runner modules run an
engine.
"""
