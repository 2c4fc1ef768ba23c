"""Sub-commands of the vcnc command line, one module each (see ``vcnc.cli``)."""
