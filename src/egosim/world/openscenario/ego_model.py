"""The ego's vehicle model built from the scenario's <Vehicle>: its bounding box, axles
and performance on the body, tyres and powertrain of egosim's ego model.

A scenario's ego is a car of stated size (Euro NCAP's test car, a catalogue's sedan):
collision timing depends on where its front is. What the file states replaces the
base model's figure; what it cannot state (tyre stiffness, inertia, drag) is the base
model's, scaled with the mass and the frontal area so that the car handles like the
base one.

- BoundingBox length, width, height and Center x: the body; the rear overhang is the
  box's reach behind the rear axle.
- Axles, FrontAxle.positionX - RearAxle.positionX: the wheelbase; the front overhang is
  the box's reach past the front axle. FrontAxle trackWidth, wheelDiameter and
  maxSteering: the track, the wheel radius and the largest front wheel angle.
- Performance maxSpeed: the governed top speed; maxDeceleration: the full-brake
  deceleration; maxAcceleration: the drive torque that gives it at the wheels.
- Vehicle mass (1.1+): the mass (none: the base model's).
"""

from __future__ import annotations

import math
from dataclasses import replace

from egosim.world.openscenario.entities import EntityDefinition
from egosim.world.vehicle.catalogue import VehicleModel


class UnusableFiguresError(ValueError):
    """The scenario's figures do not make a car (the message says which)."""


def scenario_ego_model(definition: EntityDefinition, base: VehicleModel) -> VehicleModel:
    """`base` with the body, axles and performance `definition` states.

    Without <Axles> the base model's wheelbase is kept and placed in the box from its
    rear axle; UnusableFiguresError when the figures cannot describe a car (a
    wheelbase longer than the box, a non-positive size)."""
    length, width, height = definition.length, definition.width, definition.height
    if not all(math.isfinite(v) and v > 0.0 for v in (length, width, height)):
        raise UnusableFiguresError(f"a bounding box of {length} x {width} x {height} m")
    rear_overhang = length / 2.0 - definition.centre[0]
    figures = definition.figures
    if figures is not None:
        wheelbase = figures.front_axle_x - figures.rear_axle_x
        rear_overhang += figures.rear_axle_x
    else:
        wheelbase = base.wheelbase
    front_overhang = length - wheelbase - rear_overhang
    if not (wheelbase > 0.0 and rear_overhang >= 0.0 and front_overhang >= 0.0):
        raise UnusableFiguresError(
            f"axles {wheelbase:.3f} m apart do not fit a {length:.3f} m box "
            f"({rear_overhang:.3f} m behind the rear axle)"
        )
    mass = base.mass
    if figures is not None and figures.mass is not None and figures.mass > 0.0:
        mass = figures.mass
    mass_ratio = mass / base.mass
    area_ratio = (width * height) / (base.width * base.height)
    # The base's axle-load split and yaw dynamic index carry over to the new wheelbase.
    rear_share = base.cg_to_rear_axle / base.wheelbase
    cg_to_rear = rear_share * wheelbase
    cg_to_front = wheelbase - cg_to_rear
    yaw_index = base.yaw_inertia / (base.mass * base.cg_to_front_axle * base.cg_to_rear_axle)
    model = replace(
        base,
        name=definition.model,
        length=length,
        width=width,
        height=height,
        wheelbase=wheelbase,
        front_overhang=front_overhang,
        rear_overhang=rear_overhang,
        mass=mass,
        yaw_inertia=yaw_index * mass * cg_to_front * cg_to_rear,
        cg_to_front_axle=cg_to_front,
        cg_to_rear_axle=cg_to_rear,
        cg_height=base.cg_height * height / base.height,
        cornering_stiffness_front=base.cornering_stiffness_front * mass_ratio,
        cornering_stiffness_rear=base.cornering_stiffness_rear * mass_ratio,
        max_power=base.max_power * mass_ratio,
        drag_area=base.drag_area * area_ratio,
    )
    if figures is not None:
        if figures.track_width > 0.0:
            model = replace(model, track_width=figures.track_width)
        if figures.wheel_diameter > 0.0:
            torque_per_radius = model.max_drive_torque / model.wheel_radius
            model = replace(
                model,
                wheel_radius=figures.wheel_diameter / 2.0,
                max_drive_torque=torque_per_radius * figures.wheel_diameter / 2.0,
            )
        if 0.0 < figures.max_steering < math.pi / 2.0:
            model = replace(model, max_steer_front=figures.max_steering)
    if math.isfinite(definition.max_speed) and definition.max_speed > 0.0:
        model = replace(model, max_speed=definition.max_speed)
    if math.isfinite(definition.max_deceleration) and definition.max_deceleration > 0.0:
        model = replace(model, max_brake_decel=definition.max_deceleration)
    if math.isfinite(definition.max_acceleration) and definition.max_acceleration > 0.0:
        model = replace(
            model, max_drive_torque=mass * definition.max_acceleration * model.wheel_radius
        )
    return model
