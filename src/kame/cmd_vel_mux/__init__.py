"""yocs_cmd_vel_mux: several velocity commanders, one base; the highest-priority commander that
is still talking drives. `selection` is the rule (pure), `node` the ROS node."""
