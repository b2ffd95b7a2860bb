"""dynamic_reconfigure in kame: the .cfg generator and the Config modules it makes with no build step."""
