"""interpolators package."""
