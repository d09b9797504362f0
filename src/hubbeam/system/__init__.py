"""The hub-beam system: beam meshes, hub kinematics, constraints, loads and assembly."""
