"""The files the project reads and writes beside bags and pattern libraries (no rclpy).

- :mod:`.config`: THE place config files are found (:func:`~.config.config_file`: the source
  tree's ``config/``, else the installed package's ``share/backlash_monitor/config/``) and the
  one-line messages for what is wrong in one (where YAML broke, the nearest valid key).
- :mod:`.outputs`: outputs that never destroy data (no writing over an input or, without
  ``--overwrite``, over an existing file; written under a temporary name, renamed when complete).
"""
