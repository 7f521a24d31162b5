"""Tools for teaching a class with camlab: graded assignments and lecture mode.

* :mod:`camlab.classroom.lessons` finds a lesson notebook by number or name;
* :mod:`camlab.classroom.assignments` turns lessons into an nbgrader course directory
  (``camlab assignments DEST [LESSON ...]``);
* :mod:`camlab.classroom.present` serves one lesson's demos without code through Voila
  (``camlab present 07``).

See ``docs/teaching.md`` for Binder, a JupyterHub for a class, and sizing.
"""
