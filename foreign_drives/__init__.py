"""foreign_drives: a second, independent generator of drive recordings (docs/foreign_drives.md)."""
