"""Backlash-width classifier cores (no rclpy): the paper's counter-propagation network, the improved
shape mode, fusion of consecutive onset events and the versioned pattern library.

See docs/classifier.md.
"""
