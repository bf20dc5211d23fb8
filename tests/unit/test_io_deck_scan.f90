!> Deck scanning and checking without a run: value texts of the keys, the
!> type and finiteness check, the did-you-mean guess, the restart comparison
!> of two decks, the key tables of the deck groups, and the ETA from the
!> recent rate.
program test_io_deck_scan
  use core_kinds, only: rk
  use core_status, only: status_t
  use io_deck_scan, only: deck_scan, group_instance_t, value_problem, edit_distance, &
      closest_name, LINE_LEN
  use io_deck, only: deck_restart_check, deck_known_keys, deck_group_keys, &
      DECK_GROUPS
  use core_keys, only: key_t
  use solver_eta, only: eta_t
  use check, only: check_true, check_close, check_summary
  implicit none
  character(len=LINE_LEN), allocatable :: lines(:)
  type(group_instance_t), allocatable :: groups(:)
  type(status_t) :: status
  type(eta_t) :: eta
  integer :: ngroup, g, k
  type(key_t), allocatable :: keys(:)
  logical :: tables_ok
  character(len=*), parameter :: NL = achar(10)
  character(len=:), allocatable :: base

  ! Value texts: comments and blanks dropped, blanks between items a comma,
  ! multi-line arrays joined, quoted text kept as it is.
  lines = [character(len=LINE_LEN) :: &
      "&mesh x = 0.0,  1.0 ! the ends", &
      "   nx = 10  y = 0.0 0.5", &
      "   1.0, name = 'a, b = c' /"]
  call deck_scan(lines, groups, ngroup, status)
  call check_true('one group, no problem', ngroup == 1 .and. status%ok())
  call check_true('four keys', groups(1)%nkey == 4)
  call check_true('x value', groups(1)%value(1) == '0.0,1.0')
  call check_true('nx value', groups(1)%value(2) == '10')
  call check_true('y value over two lines', groups(1)%value(3) == '0.0,0.5,1.0')
  call check_true('quoted value kept', groups(1)%value(4) == '''a, b = c''')

  ! Types and finiteness.
  call check_true('real ok', value_problem('1.0,-2,3.5d-3,.5,2*1e3', 'r') == '')
  call check_true('real overflow', index(value_problem('1.0e400', 'r'), 'not a finite') > 0)
  call check_true('real inf', index(value_problem('0.0,-Inf', 'r'), '''-Inf'' is not a finite') > 0)
  call check_true('real largest', value_problem('1.7976931348623157e308,179.7e306', 'r') == '')
  call check_true('real just above', index(value_problem('1.7976931348623158e308', 'r'), &
      'not a finite') > 0)
  call check_true('real 1e309', index(value_problem('0.001e312', 'r'), 'not a finite') > 0)
  call check_true('real tiny', value_problem('1e-400,0.0e999,-0.0', 'r') == '')
  call check_true('real nan', index(value_problem('NaN', 'r'), 'not a finite') > 0)
  call check_true('real text', index(value_problem('''abc''', 'r'), '''abc'' is not a real') > 0)
  call check_true('real 1.4.2', index(value_problem('1.4.2', 'r'), 'not a real') > 0)
  call check_true('integer ok', value_problem('10,0,3*2', 'i') == '')
  call check_true('integer real', index(value_problem('1.5', 'i'), 'not an integer') > 0)
  call check_true('integer range', index(value_problem('99999999999', 'i'), 'range') > 0)
  call check_true('logical ok', value_problem('.true.,F,.f.,T', 'l') == '')
  call check_true('logical number', index(value_problem('2', 'l'), 'not a logical') > 0)
  call check_true('string ok', value_problem('''box'',"a b"', 'c') == '')
  call check_true('string unquoted', index(value_problem('box', 'c'), 'in quotes') > 0)
  call check_true('null values', value_problem(',,1.0', 'r') == '')

  ! Every group's key table: names given once (and not cut short by the
  ! table's name length), a type, a default and a meaning for each, no '|'
  ! (the --keys field separator); the names the checks use are the table's.
  do g = 1, size(DECK_GROUPS)
    keys = deck_group_keys(trim(DECK_GROUPS(g)))
    tables_ok = size(keys) > 0 .and. all(deck_known_keys(trim(DECK_GROUPS(g))) == keys%name)
    do k = 1, size(keys)
      tables_ok = tables_ok .and. count(keys%name == keys(k)%name) == 1 .and. &
          len_trim(keys(k)%name) < len(keys(k)%name) .and. &
          index('rilc', keys(k)%type) > 0 .and. len_trim(keys(k)%default) > 0 .and. &
          len_trim(keys(k)%meaning) > 0 .and. index(keys(k)%default, '|') == 0 .and. &
          index(keys(k)%units, '|') == 0 .and. index(keys(k)%meaning, '|') == 0
    end do
    call check_true('key table of &'//trim(DECK_GROUPS(g)), tables_ok)
  end do
  call check_true('no keys for an unknown group', size(deck_group_keys('colour')) == 0)

  ! Did you mean.
  call check_true('distance tend t_end', edit_distance('tend', 't_end') == 1)
  call check_true('distance gama gamma', edit_distance('gama', 'gamma') == 1)
  call check_true('guess t_end', closest_name('tend', deck_known_keys('control')) == 't_end')
  call check_true('guess max_cycles', &
      closest_name('max_cycle', deck_known_keys('control')) == 'max_cycles')
  call check_true('no guess for colour', closest_name('colour', deck_known_keys('control')) == '')
  call check_true('guess control', closest_name('contorl', DECK_GROUPS) == 'control')

  ! Restart comparison: comments, blanks, key order and &control / &output
  ! may change; anything else is named.
  base = "&control t_end = 1.0, cfl = 0.5 /"//NL//"&mesh x = 0.0, 1.0, nx = 10 /"//NL// &
      "&material name = 'gas', eos = 'ideal_gas', gamma = 1.4 /"//NL// &
      "&output dump_cycles = 10 /"//NL
  call status%clear()
  call deck_restart_check(base, base, status)
  call check_true('same deck passes', status%ok())
  call deck_restart_check(base, "! comment"//NL//"&control t_end = 2.0 /"//NL// &
      "&mesh  nx = 10,"//NL//"  x = 0.0 1.0 ! ends"//NL//"/"//NL// &
      "&material gamma=1.4, name='gas', eos='ideal_gas' /"//NL//"&output /"//NL, status)
  call check_true('reformatted deck, new t_end and &output pass', status%ok())
  call deck_restart_check(base, "&control t_end = 1.0, cfl = 0.5 /"//NL// &
      "&mesh x = 0.0, 1.0, nx = 12 /"//NL// &
      "&material name = 'gas', eos = 'ideal_gas', gamma = 1.6 /"//NL// &
      "&output dump_cycles = 10 /"//NL, status)
  call check_true('two changes found', status%count == 2)
  if (status%count == 2) then
    call check_true('nx named', index(status%messages(1), '&mesh: nx: changed') == 1)
    call check_true('gamma named', index(status%messages(2), '&material(1): gamma: changed') == 1)
  end if
  call status%clear()
  call deck_restart_check(base, base//"&material name = 'air', eos = 'ideal_gas', gamma = 1.4 /", &
      status)
  call check_true('an added &material found', status%count == 1)
  call status%clear()
  call deck_restart_check(base, "&control t_end = 1.0 /"//NL//"&mesh x = 0.0, 1.0, nx = 10 /"// &
      NL//"&material name = 'gas', eos = 'ideal_gas' /"//NL//"&hydro q_linear = 0.2 /", status)
  call check_true('removed gamma and added &hydro found', status%count == 2)

  ! ETA from the recent rate: the newest five intervals only.
  call check_true('no eta from one sample', eta%seconds_left(1.0_rk) < 0.0_rk)
  call eta%add(0.0_rk, 0.0_rk)
  call eta%add(100.0_rk, 0.1_rk) ! slow start: 1e-3 per second
  do g = 1, 5
    call eta%add(100.0_rk + g, 0.1_rk + 0.01_rk * g) ! then 1e-2 per second
  end do
  call check_close('eta at the recent rate', eta%seconds_left(1.0_rk), (1.0_rk - 0.15_rk) / &
      0.01_rk, 1.0e-12_rk)

  call check_summary()
end program test_io_deck_scan
