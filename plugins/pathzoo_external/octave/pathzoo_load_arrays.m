## -*- texinfo -*-
## @deftypefn {} {@var{problem} =} pathzoo_load_arrays (@var{problem})
## Replace the arrays pathzoo wrote to .npy files (large maps) by their values.
##
## pathzoo writes an array of more than 65536 cells to a file and puts the
## file's path in its field; the function then sees a matrix either way.
## @end deftypefn

function problem = pathzoo_load_arrays (problem)
  for field = {"occupancy", "elevation"}
    if (isfield (problem, field{1}) && ischar (problem.(field{1})))
      problem.(field{1}) = pathzoo_read_npy (problem.(field{1}));
    endif
  endfor
  if (isfield (problem, "rules") && ischar (problem.rules.soil_strength))
    problem.rules.soil_strength = pathzoo_read_npy (problem.rules.soil_strength);
  endif
endfunction
