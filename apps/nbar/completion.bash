# bash completion for nbar: installed as /usr/share/bash-completion/completions/nbar.
# The commands and each command's options are read from the program's own --help when asked,
# so they are never out of step with the program; everything else completes as a file name.
_nbar() {
  local current="${COMP_WORDS[COMP_CWORD]}"
  local program="${COMP_WORDS[0]}"
  local command="" word previous=""
  # The command is the first word that is neither an option nor --lang's value (nbar --lang es check).
  for word in "${COMP_WORDS[@]:1:COMP_CWORD-1}"; do
    case "$word" in -*) ;; *) [ "$previous" != "--lang" ] && { command="$word"; break; } ;; esac
    previous="$word"
  done
  if [ "${COMP_WORDS[COMP_CWORD-1]}" = "--lang" ]; then
    COMPREPLY=($(compgen -W "en es" -- "$current"))
    return
  fi
  if [ -z "$command" ]; then
    local commands
    commands="$("$program" --help 2>/dev/null | awk '/^Subcommands:/{listing = 1; next} listing && /^  [a-z]/{print $1} listing && /^$/{exit}')"
    COMPREPLY=($(compgen -W "$commands --help --version --lang" -- "$current"))
    return
  fi
  if [[ "$current" == -* ]]; then
    local options
    options="$("$program" "$command" --help 2>/dev/null | grep -o -- '--[a-z][a-z0-9-]*' | sort -u)"
    COMPREPLY=($(compgen -W "$options" -- "$current"))
    return
  fi
  COMPREPLY=($(compgen -f -- "$current"))
  compopt -o filenames 2>/dev/null
}
complete -F _nbar nbar
