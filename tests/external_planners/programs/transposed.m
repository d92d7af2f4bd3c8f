## A test planner that returns its path with one row per coordinate (x's, then y's): a wrong shape.
function [path, info] = transposed (problem, params)
  path = [problem.start(:), (problem.start(:) + problem.goal(:)) / 2, problem.goal(:)];
  info = struct ("status", "solved");
endfunction
