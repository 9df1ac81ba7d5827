"""Reports: text tables and Matplotlib figures of results (no printing, no backend)."""
