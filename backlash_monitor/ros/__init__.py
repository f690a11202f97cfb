"""The ROS runtime the nodes share (docs/architecture.md): not nodes themselves, no executables.

:mod:`.runtime` (init, build, spin, clean shutdown), :mod:`.lean_executor` (the executor),
:mod:`.parameters` and :mod:`.params_file` (declared, validated parameters and ``--params-file`` checks),
:mod:`.qos` (the topics' QoS profiles), :mod:`.fast_dds` (the writer profile), :mod:`.netns` (two "hosts"
on one machine), :mod:`.conversions` (messages <-> numpy), :mod:`.drive_diagnostics` (a node's
/diagnostics status) and :mod:`.model_fit_caveat` (the width's model-fit caveat, live). May import rclpy;
imported by nodes/ and commands/ only.
"""
