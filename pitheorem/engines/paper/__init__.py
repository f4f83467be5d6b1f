"""The white paper's robots as shipped files: the hinged rod (``rod``) and SUPERball (``superball``).

They are loaded and run through :func:`pitheorem.engines.load` as a
user's file is; these modules set the paper's numbers into the files and
draw the runs, and run no engine by hand.
"""
