"""The bridge's bottom storey: what the MORAI protocol is, before anything runs.

The table of every topic and service (table.py: key, MORAI name, type, direction,
default name and rate), the files that override it (network.py: MORAI's Network
Settings tab; sensor_settings.py: its `sensors:` section), the protocol's codes
(codes.py) and units (units.py: degrees and km/h, the only place they are made), the
releases it is spoken in (releases.py) and the small builders of nested standard
messages (messages.py). Nothing here imports the rest of the bridge.
"""
