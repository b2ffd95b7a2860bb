"""image_transport as kame has it: the compressed transport's codec (pure) and the republish node."""
