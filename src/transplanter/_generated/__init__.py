"""Generated modules: written by derivations/build.py, never edited by hand."""
