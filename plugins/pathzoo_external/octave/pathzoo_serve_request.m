## -*- texinfo -*-
## @deftypefn {} {@var{text} =} pathzoo_serve_request (@var{line})
## Run one request of pathzoo's Octave shim and return the reply as JSON text.
##
## The reply has three fields: @code{answer} (pathzoo's answer object),
## @code{output} (what the function printed) and @code{error} (empty, or why
## the call failed or its outputs could not be read).
## @end deftypefn

function text = pathzoo_serve_request (line)
  try
    request = jsondecode (line);
    [folder, name] = fileparts (request.file);
    if (! any (strcmp (folder, strsplit (path (), pathsep ()))))
      addpath (folder);  # slow (tens of ms): once per folder, which stays on the path
    endif
    files = dir (fullfile (folder, "*.m"));
    [~, names] = cellfun (@fileparts, {files.name}, "UniformOutput", false);
    clear (names{:});  # the folder's functions, with their persistent variables: each run starts alike
    clear -global;
    problem = pathzoo_load_arrays (request.problem);
    pathzoo_seed (problem.seed);
    n_out = nargout (name);
  catch err
    text = reply_text (struct (), "", ["could not be prepared: " err.message]);
    return;
  end_try_catch
  info = struct ();
  try
    if (n_out == 1)
      printed = evalc ("p = feval (name, problem, problem.params);");
    else
      printed = evalc ("[p, info] = feval (name, problem, problem.params);");
    endif
  catch err
    where = "";
    if (! isempty (err.stack))
      where = sprintf (" (%s, line %d)", err.stack(1).name, err.stack(1).line);
    endif
    text = reply_text (struct (), "", ["raised an error: " err.message where]);
    return;
  end_try_catch
  [answer, unreadable] = pathzoo_encode_answer (p, info);
  text = reply_text (answer, printed, unreadable);
endfunction

function text = reply_text (answer, printed, error_text)
  text = jsonencode (struct ("answer", answer, "output", printed, "error", error_text));
endfunction
