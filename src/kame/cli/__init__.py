"""kame.cli: the ros* command-line tools, one module per command."""
