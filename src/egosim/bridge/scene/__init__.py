"""The rows that serve the scene around the egos: objects, lights, scenarios, the map.

objects.py: ObjectStatusList and the collision rows; lights.py: traffic lights and
intersections; scenarios.py: ScenarioLoad by topic and service; storyboard.py: the tick
stage of an OpenSCENARIO storyboard; specs.py: MapSpec and VehicleSpec; markers.py: the
scene as RViz markers.
"""
