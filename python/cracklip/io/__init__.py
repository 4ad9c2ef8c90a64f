"""Files: scene files (TOML), results.json, CSV, ParaView (VTU) and PNG writers.
"""
