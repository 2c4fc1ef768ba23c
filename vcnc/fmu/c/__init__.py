"""C sources of the exported FMUs (package data: *.c, *.h), read by vcnc.fmu._sources."""
