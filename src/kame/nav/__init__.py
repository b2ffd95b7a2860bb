"""Navigation: amcl, move_base, gmapping algorithms (pure) and their nodes."""
