"""Python ports of the MATLAB example programs behind the white paper.

The white paper "Scaling Analysis for Rigid Body Simulations" (A. P. Sabelhaus, NTRT, 2014) was
built from a handful of MATLAB scripts in the NTRTsim repository
(``src/dev/apsabelhaus/scaling_analysis/``).  This package re-implements them in Python, one module
per MATLAB program, keeping the original numerics (forward Euler, same step, same order of floating
point operations) so that the results can be compared with the MATLAB figure files bit for bit:

``rod_hinge_dynamics``
    Right-hand side of the hinged rod (paper Eq. 1), plus the two variants that the MATLAB file
    kept commented out (longitudinal spring/damper).
``scaling_counterexample_nonlinear``
    The hinged rod under successive scalings: the paper's Figures 1-5.
``scaling_counterexample``
    Vertical spring-mass-damper (paper Section 5): linear superposition makes the naive
    "scale gravity with length" rule work.
``scaling_counterexample_projectile``
    A projectile under scaled gravity, rescaled post hoc.
``figdata``
    A small reader for MATLAB ``.fig`` files (MAT v5), used to check the ports against the
    reference figures.

Every simulation module runs on its own, ``python matlab_ports/NAME.py --outdir DIR``, and writes
its figures as PNG files (rendered with matplotlib's Agg canvas).  Quirks of the originals are kept
and marked with ``QUIRK`` comments in the code.  The package is not part of the installed
``pitheorem`` distribution; import it from the repository root::

    from matlab_ports import scaling_counterexample_nonlinear
"""
