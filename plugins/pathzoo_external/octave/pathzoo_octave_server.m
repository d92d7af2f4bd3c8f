## pathzoo's Octave shim: serve planner requests, one JSON line in, one answer line out.
##
## Started once per pathzoo worker by pathzoo_external.octave. Each request
## names a function file, a scratch folder and the problem; the answer line
## follows a marker (char 30, PATHZOO-ANSWER, char 30). Between requests the
## functions (and their persistent variables), the global variables, the
## working directory and the path are reset, so every run starts alike.

pathzoo_marker__ = char ([30, double('PATHZOO-ANSWER'), 30]);
pathzoo_home__ = pwd ();
pathzoo_path__ = path ();
fprintf (stdout, "%sready\n", pathzoo_marker__);
fflush (stdout);
while (true)
  pathzoo_line__ = fgetl (stdin);
  if (! ischar (pathzoo_line__))
    break;
  endif
  pathzoo_answer__ = pathzoo_serve_request (pathzoo_line__);
  cd (pathzoo_home__);
  path (pathzoo_path__);
  clear -f;
  clear -g;
  fprintf (stdout, "%s%s\n", pathzoo_marker__, pathzoo_answer__);
  fflush (stdout);
endwhile
