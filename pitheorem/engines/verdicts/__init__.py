"""Verdicts: a model and its scaled copy run, compared, audited, and the causes of a difference found.

``verify`` (the runs against the one-ulp yardstick), ``audit`` (every
number the engine holds against the original times its factor),
``diagnose`` (the counter-runs that show a cause), ``causes`` (the
:class:`~pitheorem.engines.Cause` record) and ``sweep`` (``verify`` at many
scale factors, on every core or a Dask cluster).  They ask a model's runner only
what :mod:`pitheorem.engines.protocols` names, and name no engine.
"""
