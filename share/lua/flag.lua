-- flag.lua: a yes/no setting given as a -v variable, where it arrives as a string or a number.
--   local flag = require("flag")
--   flag(var.one_sided, true, "one_sided")  -> true or false
-- true, 1, "1" and "true" are yes; false, 0, "0" and "false" are no; nil (not given) is
-- `default`; anything else is an error that names the variable.
return function(value, default, name)
  if value == nil then return default end
  if value == true or value == 1 or value == "1" or value == "true" then return true end
  if value == false or value == 0 or value == "0" or value == "false" then return false end
  error(string.format("variable '%s' must be true or false (or 1 or 0), got %s", name or "?", tostring(value)), 2)
end
