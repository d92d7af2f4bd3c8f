## -*- texinfo -*-
## @deftypefn {} {@var{a} =} pathzoo_read_npy (@var{file})
## Read an array pathzoo saved with numpy.save (C order; uint8, bool or float64) as a double array.
## @end deftypefn

function a = pathzoo_read_npy (file)
  [fid, msg] = fopen (file, "r", "ieee-le");
  if (fid < 0)
    error ("pathzoo_read_npy: cannot open %s: %s", file, msg);
  endif
  magic = fread (fid, 6, "uint8=>char")';
  version = fread (fid, 2, "uint8");
  if (! strcmp (magic(2:6), "NUMPY"))
    fclose (fid);
    error ("pathzoo_read_npy: %s is not an .npy file", file);
  endif
  if (version(1) == 1)
    header_length = fread (fid, 1, "uint16");
  else
    header_length = fread (fid, 1, "uint32");
  endif
  header = fread (fid, header_length, "uint8=>char")';
  descr = regexp (header, "'descr':\\s*'([^']*)'", "tokens", "once"){1};
  shape = str2num (["[" regexp(header, "'shape':\\s*\\(([^)]*)\\)", "tokens", "once"){1} "]"]);
  switch (descr)
    case {"|u1", "|b1"}
      precision = "uint8=>double";
    case "<f8"
      precision = "float64=>double";
    otherwise
      fclose (fid);
      error ("pathzoo_read_npy: %s holds %s values, not uint8, bool or float64", file, descr);
  endswitch
  data = fread (fid, prod (shape), precision);
  fclose (fid);
  a = permute (reshape (data, fliplr (shape)), numel (shape):-1:1);
endfunction
