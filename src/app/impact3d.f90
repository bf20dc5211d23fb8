!> impact3d: 3D staggered Lagrangian hydrocode with contact.
!> Usage: impact3d [--check] [--restart dump.h5 [--restart-force]] deck.nml
program impact3d
  use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
  use app_run, only: run_deck, EXIT_OK, EXIT_INPUT
  use parallel_env, only: par_init, par_finalize, par_rank
  use io_deck, only: deck_group_keys, DECK_GROUPS
  use core_keys, only: key_t, key_line
  use core_signal, only: signal_install
  use core_exit, only: process_exit
  use core_version, only: IMPACT3D_VERSION
  implicit none
  character(len=512) :: arg, deck, restart
  integer :: i, nargs, code
  logical :: check_only, ok, force

  call par_init()
  ! After MPI_Init, so that these handlers are the ones in force.
  call signal_install(ok)
  if (.not. ok) write(error_unit, '(a,i0,a)') 'rank ', par_rank(), ': impact3d: warning: '// &
      'could not install the SIGTERM/SIGUSR1/SIGUSR2 handlers: signals will kill the run'
  deck = ''
  restart = ''
  check_only = .false.
  force = .false.
  code = EXIT_OK
  nargs = command_argument_count()
  i = 0
  do while (i < nargs)
    i = i + 1
    call get_command_argument(i, arg)
    select case (trim(arg))
    case ('-h', '--help')
      if (par_rank() == 0) write(output_unit, '(a)') &
          'usage: impact3d [--check] [--restart dump.h5 [--restart-force]] deck.nml', &
          '  --version        print the version and stop', &
          '  --keys           list every deck key: group, name, type, default, units, meaning', &
          '  --materials      list the material library: parameters and sources', &
          '  --check          validate the deck and set up the mesh, run nothing', &
          '  --restart F      continue from dump F (same deck and mesh; &control and', &
          '                   &output may change)', &
          '  --restart-force  restart even though other groups of the deck changed'
      check_only = .true.
      deck = '-'
      exit
    case ('--version')
      if (par_rank() == 0) write(output_unit, '(a)') 'impact3d '//IMPACT3D_VERSION
      check_only = .true.
      deck = '-'
      exit
    case ('--restart-force')
      force = .true.
    case ('--keys')
      if (par_rank() == 0) call print_keys()
      check_only = .true.
      deck = '-'
      exit
    case ('--check')
      check_only = .true.
    case ('--materials')
      if (par_rank() == 0) call print_materials()
      check_only = .true.
      deck = '-'
      exit
    case ('--restart')
      i = i + 1
      if (i > nargs) then
        code = EXIT_INPUT
        if (par_rank() == 0) write(error_unit, '(a)') 'impact3d: --restart needs a file name'
      else
        call get_command_argument(i, restart)
      end if
    case default
      if (arg(1:1) == '-') then
        code = EXIT_INPUT
        if (par_rank() == 0) write(error_unit, '(a)') 'impact3d: unknown option '//trim(arg)
      else if (len_trim(deck) > 0) then
        code = EXIT_INPUT
        if (par_rank() == 0) write(error_unit, '(a)') 'impact3d: only one deck, please'
      else
        deck = arg
      end if
    end select
  end do
  if (code == EXIT_OK .and. len_trim(deck) == 0) then
    code = EXIT_INPUT
    if (par_rank() == 0) write(error_unit, '(a)') &
        'usage: impact3d [--check] [--restart dump.h5 [--restart-force]] deck.nml'
  end if
  if (code == EXIT_OK .and. deck /= '-') call run_deck(trim(deck), trim(restart), check_only, &
      force, code)
  call par_finalize()
  ! The exit status without 'STOP n' on standard error (the message is out).
  if (code /= EXIT_OK) call process_exit(code)
contains

  !> Every deck key, one per line: '&group | key | type | default | units |
  !> meaning' (units '-' when there are none), groups in deck order.
  subroutine print_keys()
    type(key_t), allocatable :: keys(:)
    integer :: g, k
    do g = 1, size(DECK_GROUPS)
      keys = deck_group_keys(trim(DECK_GROUPS(g)))
      do k = 1, size(keys)
        write(output_unit, '(a)') key_line(trim(DECK_GROUPS(g)), keys(k))
      end do
    end do
  end subroutine print_keys

  !> Every built-in data set: its parameters as a deck with library = name
  !> gets them (strength models with data in the set), and their source.
  subroutine print_materials()
    use material_table, only: material_t, LIBRARY_NAMES, EOS_MIE_GRUNEISEN, material_library, &
        STRENGTH_STEINBERG_GUINAN, STRENGTH_JOHNSON_COOK
    use core_kinds, only: rk
    use core_unit_checks, only: real_text => brief_text
    use material_flow_stress, only: sg_set, jc_set
    use app_summary, only: material_lines
    type(material_t) :: mat
    character(len=600), allocatable :: lines(:)
    integer :: k
    logical :: found
    write(output_unit, '(a)') 'material library (cm-g-us-mbar, K; &material library = name, '// &
        'eos = ''mie_gruneisen''; any key given overrides the library''s value):'
    do k = 1, size(LIBRARY_NAMES)
      mat = material_t()
      mat%name = LIBRARY_NAMES(k)
      mat%library = LIBRARY_NAMES(k)
      mat%eos = EOS_MIE_GRUNEISEN
      call material_library(trim(LIBRARY_NAMES(k)), mat%mg, mat%shear_modulus, &
          mat%yield_stress, found)
      write(output_unit, '(a)') '  '''//trim(LIBRARY_NAMES(k))//''':'
      lines = material_lines(mat, 'cm-g-us-mbar')
      write(output_unit, '(a)') trim(lines(1))
      ! Strength: elastic-plastic G and Y0, then the model sets the library has.
      if (mat%shear_modulus > 0.0_rk) then
        write(output_unit, '(a)') '    strength elastic_plastic: G = '// &
            real_text(mat%shear_modulus)//', Y0 = '//real_text(mat%yield_stress)
      else
        write(output_unit, '(a)') '    strength elastic_plastic: Y0 = '// &
            real_text(mat%yield_stress)//' (no G: give shear_modulus)'
      end if
      mat%sg = sg_set(trim(LIBRARY_NAMES(k)))
      if (mat%sg%g0 > 0.0_rk) then
        mat%strength = STRENGTH_STEINBERG_GUINAN
        lines = material_lines(mat, 'cm-g-us-mbar')
        write(output_unit, '(a)') trim(lines(2))
      end if
      mat%jc = jc_set(trim(LIBRARY_NAMES(k)))
      if (mat%jc%a > 0.0_rk) then
        mat%strength = STRENGTH_JOHNSON_COOK
        lines = material_lines(mat, 'cm-g-us-mbar')
        write(output_unit, '(a)') trim(lines(2))
      end if
      write(output_unit, '(a)') trim(lines(size(lines)))
    end do
  end subroutine print_materials

end program impact3d
