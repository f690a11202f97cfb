"""The live model watch's cores (docs/model_watch.md; plain numpy, no rclpy): a drive's onset events against its
model version's precomputed reference (workbench/reference.py), the alarm rule, and the evidence kept on a WARN.

- events.py: the live onset events of a stream (the workbench's event definition);
- alarm.py: when the model no longer explains the drive (measured thresholds, persistence);
- core.py: ModelWatch: the window of the last N events, evaluated after each;
- snapshot.py: the ring of the plant topics and the bag of X s before and Y s after a WARN.
"""
