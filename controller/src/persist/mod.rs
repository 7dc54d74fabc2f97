//! Persistence: what survives power-off (settings, offsets, common variables
//! #401–#600, the program store) on NOR flash.
