"""The model workbench (SPEC section 5): hold the model against a measurement, see where it fails, find the
missing physical effect, add it, watch the error fall. Plain numpy/scipy, no rclpy; docs/workbench.md.

- measurement.py: loading MCAP/CSV/NPZ recordings and checking them against a model
- model.py: versioned model YAML, --set overrides, history log; versions.py: the next version
- plant_adapter.py: the one door to the plant simulator (catalogue, shared-noise batches)
- events.py: onset segments, event averages, the model's noise ensemble
- spectral.py: the raw (not denoised) spectral shape of every onset event (the sensor roll-off's view)
- analysis.py: comparison, fit %, spread, spectra, where the residual sits
- fitting.py: candidate fits on common random numbers, uncertainty, BIC on events
- diagnose.py: the decisions; report.py: PNGs + HTML
"""
