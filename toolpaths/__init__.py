"""toolpaths package."""
