"""A module whose import fails: validation shows Python's traceback."""

raise RuntimeError("this module refuses to be imported")
