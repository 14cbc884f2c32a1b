"""MORAI's synchronous mode: the client steps the world.

sync_session.py: its state (the context's `sync`); sync_mode.py: SyncModeCmd,
WaitForTick, the commands kept for a frame and SyncModeInfo; sync_objects.py: objects
added or removed at a frame.
"""
