## A test planner that raises an error.
function [path, info] = raises (problem, params)
  path = [];
  info = struct ();
  error ("raises: the map has %d cells", numel (problem.occupancy));
endfunction
