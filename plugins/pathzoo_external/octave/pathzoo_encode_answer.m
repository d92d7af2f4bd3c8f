## -*- texinfo -*-
## @deftypefn {} {[@var{answer}, @var{problem}] =} pathzoo_encode_answer (@var{path}, @var{info})
## pathzoo's answer object from a planner function's outputs, or why they cannot be read.
##
## @var{path} must be a numeric matrix with one row per point; it is sent as a
## list of rows whatever its shape, so pathzoo can name a wrong one. Of
## @var{info}, the fields status, times, iterations, evaluations, history and
## message are sent; other fields are ignored. Without a status, a non-empty
## path means "solved" and an empty one "failed".
## @end deftypefn

function [answer, problem] = pathzoo_encode_answer (p, info)
  answer = struct ();
  problem = "";
  if (! (isnumeric (p) || islogical (p)) || ndims (p) > 2)
    problem = sprintf ("returned path as a %s of size %s, not a numeric matrix with one row per point",
                       class (p), mat2str (size (p)));
    return;
  endif
  if (! isstruct (info) || numel (info) != 1)
    problem = sprintf ("returned info as a %s, not a struct", class (info));
    return;
  endif
  answer.path = num2cell (double (p), 2);
  if (isfield (info, "status"))
    answer.status = info.status;
  elseif (isempty (p))
    answer.status = "failed";
  else
    answer.status = "solved";
  endif
  if (isfield (info, "times"))
    answer.times = num2cell (double (info.times(:)'));
  endif
  if (isfield (info, "history"))
    answer.history = num2cell (double (info.history), 2);
  endif
  for field = {"iterations", "evaluations", "message"}
    if (isfield (info, field{1}))
      answer.(field{1}) = info.(field{1});
    endif
  endfor
endfunction
