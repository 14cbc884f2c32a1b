"""The rows that serve the main ego's sensors and cameras, and the rigs behind them.

sensor_rig.py: the sensors' models, mounts and tf frames at run time (the context's
`sensors`); sensor_rows.py: /gps, /imu, /lidar3D, /radar, /tf and SensorPosControl,
with sensor_messages.py building their messages; sensor_files.py: SaveSensorData;
camera_rig.py: the renderer and the map's static scene, built once with the rig (the
context's `cameras`); camera_rows.py: the image and CameraInfo topics. The sensor
models themselves are egosim.sensors (pure).
"""
