## pathzoo's Octave shim: serve planner requests, one JSON text in, one answer line out.
##
## Started once per pathzoo worker by pathzoo_external.octave. Each request is
## a line holding its length in bytes, then that many bytes of JSON naming a
## function file, a scratch folder and the problem (a line alone is not
## enough: fgetl on a pipe returns a line only once the next byte is there).
## The answer line follows a marker (char 30, PATHZOO-ANSWER, char 30).
## Before each call the
## functions of the function file's folder (and their persistent variables)
## and the global variables are cleared, so every run starts alike; the
## folders of the function files stay on the path. The working directory is
## the server's own temporary folder (changing it costs tens of milliseconds);
## each run's scratch folder is problem.scratch.

pathzoo_marker__ = char ([30, double('PATHZOO-ANSWER'), 30]);
fprintf (stdout, "%sready\n", pathzoo_marker__);
fflush (stdout);
while (true)
  pathzoo_length__ = fgetl (stdin);
  if (! ischar (pathzoo_length__))
    break;
  endif
  pathzoo_request__ = fread (stdin, [1, str2double(pathzoo_length__)], "char=>char");
  pathzoo_answer__ = pathzoo_serve_request (pathzoo_request__);
  fprintf (stdout, "%s%s\n", pathzoo_marker__, pathzoo_answer__);
  fflush (stdout);
endwhile
